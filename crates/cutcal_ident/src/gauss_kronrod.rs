//! The 7/15-point Gauss-Kronrod rule on one panel (Kronrod 1965; nodes and weights as in
//! QUADPACK, Piessens et al. 1983, routine QK15): the nodes of `[a, b]` with their Kronrod and
//! embedded Gauss weights, and the `(K15, |K15 - G7|)` pair the adaptive rule of
//! [`crate::zone_rule`] bisects on.

/// Kronrod abscissae on [-1, 1] (non-negative half, descending), QUADPACK QK15.
const XGK: [f64; 8] = [
    0.991_455_371_120_812_6,
    0.949_107_912_342_758_5,
    0.864_864_423_359_769_1,
    0.741_531_185_599_394_4,
    0.586_087_235_467_691_1,
    0.405_845_151_377_397_2,
    0.207_784_955_007_898_5,
    0.0,
];
/// Kronrod weights matching [`XGK`], QUADPACK QK15.
const WGK: [f64; 8] = [
    0.022_935_322_010_529_22,
    0.063_092_092_629_978_55,
    0.104_790_010_322_250_2,
    0.140_653_259_715_525_9,
    0.169_004_726_639_267_9,
    0.190_350_578_064_785_4,
    0.204_432_940_075_298_9,
    0.209_482_141_084_727_8,
];
/// Gauss weights of the embedded 7-point rule, at `XGK[1], XGK[3], XGK[5], XGK[7]`, QUADPACK QK15.
const WG: [f64; 4] =
    [0.129_484_966_168_869_7, 0.279_705_391_489_276_7, 0.381_830_050_505_118_9, 0.417_959_183_673_469_4];

/// The 15 Kronrod nodes of `[a, b]` with their Kronrod and (embedded) Gauss weights.
pub(crate) fn panel_nodes(a: f64, b: f64) -> [(f64, f64, f64); 15] {
    let c = 0.5 * (a + b);
    let hw = 0.5 * (b - a);
    let mut out = [(0.0, 0.0, 0.0); 15];
    let mut k = 0;
    for (j, (&x, &w)) in XGK.iter().zip(&WGK).enumerate() {
        let wg = if j % 2 == 1 { WG[j / 2] } else { 0.0 };
        if x == 0.0 {
            out[k] = (c, w * hw, wg * hw);
            k += 1;
        } else {
            out[k] = (c - hw * x, w * hw, wg * hw);
            out[k + 1] = (c + hw * x, w * hw, wg * hw);
            k += 2;
        }
    }
    out
}

/// `(K15, |K15 - G7|)` of `f` over `[a, b]`.
///
/// **Source:** Gauss-Kronrod 7/15 rule (Kronrod 1965; QUADPACK QK15, Piessens et al. 1983).
pub fn gauss_kronrod_15(f: impl Fn(f64) -> f64, a: f64, b: f64) -> (f64, f64) {
    let (mut k, mut g) = (0.0, 0.0);
    for (x, wk, wg) in panel_nodes(a, b) {
        let v = f(x);
        k += wk * v;
        g += wg * v;
    }
    (k, (k - g).abs())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kronrod_rule_is_exact_to_degree_22_and_gauss_to_13() {
        // Independent check: int_{-1}^{1} x^k dx = 2/(k+1) for even k, 0 for odd k.
        for k in 0..=23 {
            let exact = if k % 2 == 0 { 2.0 / (k as f64 + 1.0) } else { 0.0 };
            let nodes = panel_nodes(-1.0, 1.0);
            let kr: f64 = nodes.iter().map(|n| n.1 * n.0.powi(k)).sum();
            let ga: f64 = nodes.iter().map(|n| n.2 * n.0.powi(k)).sum();
            if k <= 22 {
                assert!((kr - exact).abs() < 1e-14, "K15 degree {k}: {kr} vs {exact}");
            }
            if k <= 13 {
                assert!((ga - exact).abs() < 1e-14, "G7 degree {k}: {ga} vs {exact}");
            }
        }
        // G7 is not exact at degree 14 (it is a 7-point Gauss rule): the error estimate is live.
        let nodes = panel_nodes(-1.0, 1.0);
        let ga: f64 = nodes.iter().map(|n| n.2 * n.0.powi(14)).sum();
        assert!((ga - 2.0 / 15.0).abs() > 1e-6);
    }

    #[test]
    fn gauss_kronrod_integrates_a_smooth_function() {
        // int_0^1 exp(x) dx = e - 1.
        let (k, e) = gauss_kronrod_15(f64::exp, 0.0, 1.0);
        assert!((k - (std::f64::consts::E - 1.0)).abs() < 1e-15);
        assert!(e < 1e-12);
    }
}
