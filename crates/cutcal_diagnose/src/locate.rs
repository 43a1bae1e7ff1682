//! Locate the mismatch (design note Sec 3.2): per output, the mean log residual with its z-test at
//! the noise level, and the strongest trend against 1/h, ln V and run order by ordinary least
//! squares.

use cutcal_model::CuttingTest;

use crate::fit::{output, Obs, OUTPUTS};
use crate::report::*;
use crate::simulator::Prediction;
use crate::stats;

/// Locates the mismatch per output: bias and the strongest covariate trend of the relative residual.
pub(crate) fn locate(
    tests: &[CuttingTest],
    obs: &[Obs],
    preds: &[Prediction],
    noise: &[f64; crate::fit::NOUT],
) -> Vec<Mismatch> {
    let mut out = Vec::new();
    for j in 0..crate::fit::NOUT {
        let rows: Vec<&Obs> = obs.iter().filter(|o| o.output == j).collect();
        if rows.is_empty() {
            continue;
        }
        let r: Vec<f64> = rows.iter().map(|o| (o.value / output(&preds[o.test], j)).ln()).collect();
        let nj = r.len() as f64;
        let mean = r.iter().sum::<f64>() / nj;
        let bias_pct = 100.0 * rows.iter().map(|o| o.value / output(&preds[o.test], j) - 1.0).sum::<f64>() / nj;
        let z = mean / (noise[j] / nj.sqrt());
        let p_bias = 2.0 * stats::normal_sf(z.abs());
        let mut trends: Vec<(String, f64, f64)> = Vec::new();
        if rows.len() >= 4 {
            let covs: Vec<(&str, Vec<Option<f64>>)> = vec![
                ("1/h", rows.iter().map(|o| Some(1e-3 / tests[o.test].uncut_chip_thickness_m)).collect()),
                ("ln V", rows.iter().map(|o| Some((tests[o.test].speed_m_per_s * 60.0).ln())).collect()),
                ("shear-zone temperature", rows.iter().map(|o| preds[o.test].t_ab_c).collect()),
                ("test order", rows.iter().map(|o| tests[o.test].order.map(f64::from)).collect()),
            ];
            for (name, c) in covs {
                if c.iter().any(Option::is_none) {
                    continue;
                }
                let x: Vec<f64> = c.into_iter().flatten().collect();
                if let Some((slope, p)) = ols_slope(&x, &r) {
                    trends.push((name.to_string(), slope, p));
                }
            }
        }
        let m = trends.len().max(1) as f64;
        let best = trends.iter().min_by(|a, b| a.2.total_cmp(&b.2));
        let (trend, p_trend) = match best {
            Some((name, slope, p)) if (p * m).min(1.0) < 0.05 => {
                let dir = if *slope > 0.0 { "rises" } else { "falls" };
                (format!("{dir} with {name} (p = {:.1e})", (p * m).min(1.0)), (p * m).min(1.0))
            }
            _ => ("none".to_string(), 1.0),
        };
        let tests_out: Vec<String> = rows
            .iter()
            .zip(&r)
            .filter(|(_, v)| v.abs() > 2.0 * noise[j])
            .map(|(o, _)| tests[o.test].id.clone())
            .collect();
        out.push(Mismatch {
            output: OUTPUTS[j].into(),
            bias_pct,
            trend,
            p_value: p_bias.min(p_trend),
            tests: tests_out,
        });
    }
    out
}

/// OLS slope of `y` on `x` with an intercept and its two-sided p-value; `None` without spread.
pub(crate) fn ols_slope(x: &[f64], y: &[f64]) -> Option<(f64, f64)> {
    let n = x.len() as f64;
    let mx = x.iter().sum::<f64>() / n;
    let my = y.iter().sum::<f64>() / n;
    let sxx: f64 = x.iter().map(|v| (v - mx).powi(2)).sum();
    if sxx <= 1e-12 * (1.0 + mx * mx) * n {
        return None;
    }
    let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let b = sxy / sxx;
    let rss: f64 = x.iter().zip(y).map(|(a, c)| (c - my - b * (a - mx)).powi(2)).sum();
    let df = n - 2.0;
    if df < 1.0 {
        return None;
    }
    let se = (rss / df / sxx).sqrt();
    let t = if se > 0.0 { b / se } else { f64::INFINITY };
    Some((b, stats::t_two_sided_p(t, df)))
}
