//! The F-test of a mechanism's refit and the parameter counts it rests on (design note Sec 3.4):
//! which parameters sit on a bound under the null (the chi-bar-square mixture of Self & Liang 1987),
//! which only shape a mechanism (no numerator degree of freedom), which are chosen on a grid
//! (counted in the AICc), and the cosine of two fitted corrections (the ambiguity rule).

use crate::context::Context;
use crate::mechanism::{info, MechanismId};
use crate::stats;

/// How many of a mechanism's fitted parameters have their off value on a bound of their range
/// (edge radius, wear land, size-effect length, built-up-edge rake shift: 0 at the lower bound;
/// friction: m_f0 = 1 at the upper and p_v = 0 at the lower bound). Under the null such a parameter
/// can only move one way, so the likelihood-ratio statistic is a chi-bar-square mixture rather than
/// chi-square(d) (Self & Liang 1987). The built-up-edge onset is chosen on a grid, not fitted.
pub(crate) fn boundary_params(id: MechanismId) -> usize {
    let inf = info(id);
    let fitted = if id == MechanismId::BuiltUpEdge { 1 } else { inf.params.len() };
    inf.params[..fitted - shape_params(id)].iter().filter(|p| p.off <= p.lower || p.off >= p.upper).count()
}

/// Fitted parameters that only shape a mechanism and have no effect when its strength is off (the
/// size effect's `w_chip` and `w_ref` at l = 0, the edge's `w_rake` at r_e = 0, the wear's running-in share
/// `w_0` at VB = 0): they are last in its list, add
/// no numerator degree of freedom to its F-test (unidentified under the null, so the test is on the
/// strength; the calibrated null refits them in every replicate, which accounts for their
/// selection), and count in the AICc and the residual degrees of freedom as any fitted parameter
/// does.
pub(crate) fn shape_params(id: MechanismId) -> usize {
    match id {
        MechanismId::SizeEffect => 2,
        MechanismId::EdgePloughing | MechanismId::FlankWear => 1,
        _ => 0,
    }
}

/// Numerator degrees of freedom of mechanism `id`'s F-test when the fit gained `added` parameters
/// with it: its shape parameters are not tested ([`shape_params`]).
pub(crate) fn tested_df(id: MechanismId, added: usize) -> usize {
    added.saturating_sub(shape_params(id))
}

/// Parameters of a mechanism chosen on a grid rather than fitted (the built-up-edge onset, its
/// floor when the gate is a band, `Context::bue_floor`, the speed when it was chosen as the
/// gate's coordinate over the interface temperature, `Context::bue_by_speed`: the temperature is
/// the edge's physical gate, the speed the alternative that has to pay; and the sharp gate's width
/// when it was chosen over the default, `Context::bue_sharp`): they count in the AICc as
/// any fitted parameter does (Burnham & Anderson 2002, Sec 2.2: K is every estimated parameter), so
/// that a mechanism with a grid-chosen gate has no advantage over one whose second parameter is
/// fitted.
pub(crate) fn grid_chosen(id: MechanismId, ctx: &Context) -> usize {
    if id == MechanismId::BuiltUpEdge {
        1 + usize::from(ctx.bue_floor > 0.0) + usize::from(ctx.bue_by_speed) + usize::from(ctx.bue_sharp_gate())
    } else {
        0
    }
}

/// Whether a refit is significant: its F-test below the round's level `alpha` and its AICc below
/// the current model's (`daicc < 0`). The F-test asks whether the data demand the mechanism; the
/// AICc, which ranks rival explanations and also counts the nuisance's prior penalty and the
/// grid-chosen gates, asks whether the model with it is better supported than the model without
/// it (Burnham & Anderson 2002, Sec 2.6). A claim that the ranking criterion itself places below
/// the current model is not made. The calibrated null (`crate::null`) sets `alpha` on the F-test
/// alone, so this condition only removes claims and the family-wise level still bounds the
/// false-positive rate.
pub(crate) fn supported(p: f64, alpha: f64, daicc: f64) -> bool {
    p.is_finite() && p < alpha && daicc < 0.0
}

/// The reason a refit is not significant in the sense of [`supported`].
pub(crate) fn unsupported_reason(p: f64, alpha: f64, daicc: f64) -> String {
    if p < alpha {
        format!(
            "its F-test passes (p = {p:.2e} < {alpha:.4}), but its AICc is no better than the model's without it \
             (dAICc {daicc:+.1}): the parameters it adds are not supported"
        )
    } else {
        format!("not significant (p = {p:.2e} >= {alpha:.4})")
    }
}

/// Binomial coefficient for the small counts of the mixture weights.
fn choose(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// F-test p-value of a nested least-squares comparison with `boundary` of its `d` new parameters
/// off on a bound of their range.
///
/// With `X = (rss0 - rss1) / s2`, the statistic of `d` parameters of which `b` sit on a bound under
/// the null is the mixture `sum_j C(b, j) 2^-b chi2(d - b + j)` (Self & Liang 1987, Theorem 3, for
/// information that is block-diagonal between the parameters; chi2(0) is a point mass at 0), each
/// component taken as its F analogue `F(q, df2)` at `X / q`. One one-sided parameter (`d = b = 1`)
/// gives the familiar halving of the two-sided p-value; `b = 0` the plain F-test.
///
/// The residuals are in units of the noise model, so the residual variance is never taken below 1:
/// a fit closer than the stated measurement scatter does not make a smaller improvement
/// significant (the test is then the known-variance one, with F(d, df2) as its conservative
/// reference). Without the floor, noise-free or over-smoothed recordings let a 0.4 % systematic
/// difference pass as physics.
pub(crate) fn f_test(rss0: f64, rss1: f64, d: usize, n: usize, k1: usize, boundary: usize) -> f64 {
    if d == 0 || n <= k1 || rss1 <= 0.0 {
        return f64::NAN;
    }
    let df2 = (n - k1) as f64;
    let x = (rss0 - rss1).max(0.0) / (rss1 / df2).max(1.0);
    let b = boundary.min(d);
    let w = 0.5f64.powi(b as i32);
    (0..=b)
        .map(|j| {
            let q = d - b + j;
            if q == 0 {
                0.0
            } else {
                choose(b, j) * w * stats::f_sf(x / q as f64, q as f64, df2)
            }
        })
        .sum()
}

pub(crate) fn cosine(a: &[f64], b: &[f64]) -> f64 {
    let (mut ab, mut aa, mut bb) = (0.0, 0.0, 0.0);
    for (x, y) in a.iter().zip(b) {
        ab += x * y;
        aa += x * x;
        bb += y * y;
    }
    if aa <= 0.0 || bb <= 0.0 {
        0.0
    } else {
        (ab / (aa * bb).sqrt()).abs()
    }
}

#[cfg(test)]
mod tests {
    use super::{boundary_params, f_test, shape_params, supported, unsupported_reason};
    use crate::mechanism::MechanismId;

    #[test]
    fn boundary_mixture_matches_the_chi_bar_square_by_hand() {
        // Large df2 (F(q, df2) q -> chi2(q)) and X = rss0 - rss1 = 6 (rss1 / df2 < 1, so s2 = 1).
        // Two parameters, both off on a bound (friction): 1/4 chi2(0) + 1/2 chi2(1) + 1/4 chi2(2).
        // P(chi2(1) > 6) = erfc(sqrt(3)) = 0.014306, P(chi2(2) > 6) = exp(-3) = 0.049787, so
        // p = 0.5 0.014306 + 0.25 0.049787 = 0.019600.
        let p = f_test(6.5, 0.5, 2, 1_000_002, 2, 2);
        assert!((p - 0.019600).abs() < 2e-4, "{p}");
        // One of two on a bound: 1/2 chi2(1) + 1/2 chi2(2) = 0.032047.
        let p = f_test(6.5, 0.5, 2, 1_000_002, 2, 1);
        assert!((p - 0.032047).abs() < 2e-4, "{p}");
        // None on a bound: the plain chi2(2) tail.
        let p = f_test(6.5, 0.5, 2, 1_000_002, 2, 0);
        assert!((p - 0.049787).abs() < 2e-4, "{p}");
        // The mechanisms' own counts: friction has both, the edge its one, softening none; the
        // built-up edge counts only its fitted rake shift (the onset is chosen on a grid).
        assert_eq!(boundary_params(MechanismId::ToolChipFriction), 2);
        assert_eq!(boundary_params(MechanismId::EdgePloughing), 1);
        assert_eq!(boundary_params(MechanismId::ThermalSoftening), 0);
        assert_eq!(boundary_params(MechanismId::BuiltUpEdge), 1);
        assert_eq!(boundary_params(MechanismId::ForceCrosstalk), 0);
        // The size effect's strength l sits at its bound; its shapes w_chip and w_ref are not tested.
        assert_eq!(boundary_params(MechanismId::SizeEffect), 1);
        assert_eq!(shape_params(MechanismId::SizeEffect), 2);
        assert_eq!(shape_params(MechanismId::FlankWear), 1);
    }

    #[test]
    fn f_test_never_takes_the_residual_variance_below_the_noise() {
        // n = 31, k1 = 1: df2 = 30. A fit far closer than the noise (rss1 = 0.01) improving the
        // RSS by 3.0 noise units: the variance is floored at 1, so F = 3.0 and, as F(1, 30) = t(30)^2,
        // p is the two-sided t(30) tail at sqrt(3) = 1.732, between the table's 0.10 (t = 1.697)
        // and 0.05 (t = 2.042), about 0.094. Without the floor F would be 9000 and p ~ 1e-35.
        let p = f_test(3.01, 0.01, 1, 31, 1, 0);
        assert!(p > 0.09 && p < 0.10, "{p}");
        // At or above the noise the data's own variance is used: rss1 = 60 on 30 df gives s2 = 2,
        // F = 30 / 2 = 15; one-sided halving for a one-sided parameter.
        let two = f_test(90.0, 60.0, 1, 31, 1, 0);
        let one = f_test(90.0, 60.0, 1, 31, 1, 1);
        assert!((one - 0.5 * two).abs() < 1e-15 && two < 1e-3 && two > 1e-4, "{two}");
    }

    #[test]
    fn a_claim_needs_its_f_test_and_an_aicc_below_the_model_without_it() {
        assert!(supported(1e-4, 0.01, -0.5));
        // Significant by its F-test, but the AICc ranks the model without it higher (a size effect
        // with five conditions on a gain decoy: dAICc +15.8).
        assert!(!supported(1e-4, 0.01, 15.8));
        assert!(!supported(1e-4, 0.01, 0.0));
        assert!(!supported(0.02, 0.01, -20.0));
        assert!(!supported(f64::NAN, 0.01, -20.0));
        let r = unsupported_reason(1e-4, 0.01, 15.8);
        assert!(r.starts_with("its F-test passes (p = 1.00e-4 < 0.0100)") && r.contains("dAICc +15.8"), "{r}");
        assert_eq!(unsupported_reason(0.02, 0.01, -20.0), "not significant (p = 2.00e-2 >= 0.0100)");
    }
}
