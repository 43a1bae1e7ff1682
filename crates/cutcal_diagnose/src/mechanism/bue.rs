//! The built-up edge's gate (design note M9; Trent & Wright 2000): the smooth indicator on its gate
//! coordinate (the interface temperature, or the speed) and the candidate onsets the fitter chooses
//! from.

use cutcal_model::CuttingTest;

use crate::context::Context;

/// Smooth indicator of the built-up edge on its gate coordinate (interface temperature, degC, or
/// speed, m/min; `Context::bue_coordinate`): 1 well below the onset, 0 well above.
#[must_use]
pub fn bue_indicator(coordinate: f64, onset: f64) -> f64 {
    // Logistic in the log of the coordinate with a width of 10 % of the onset.
    1.0 / (1.0 + ((coordinate.max(1e-9) / onset.max(1e-9)).ln() / 0.1).exp())
}

/// Candidate built-up-edge onsets on the gate coordinate: geometric midpoints between its distinct
/// values that leave at least a third of them (and at least two) out of the BUE regime; at most 8,
/// evenly spread over the ranks. An edge over nearly every condition is a uniform rake change, which
/// friction or softening explains as well: the onset is identified only with conditions on both
/// sides (with two above it, friction and softening datasets were named `built_up_edge`).
#[must_use]
pub fn bue_onsets(tests: &[CuttingTest], ctx: &Context) -> Vec<f64> {
    let mut v: Vec<f64> = (0..tests.len()).map(|i| ctx.bue_coordinate(tests, i)).filter(|x| *x > 0.0).collect();
    v.sort_by(f64::total_cmp);
    v.dedup_by(|a, b| (*a - *b).abs() <= 1e-3 * b.abs());
    if v.len() < 2 {
        return Vec::new();
    }
    let above = 2.max(v.len().div_ceil(3));
    let all: Vec<f64> = v.windows(2).map(|w| (w[0] * w[1]).sqrt()).take(v.len().saturating_sub(above).max(1)).collect();
    if all.len() <= 8 {
        return all;
    }
    (0..8).map(|k| all[k * (all.len() - 1) / 7]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bue_onsets_leave_a_third_of_the_gate_values_above() {
        // Nine interface temperatures 400, 450, ..., 800 degC: a third (3) must stay above the
        // onset, so the candidates are the 6 midpoints below the seventh value, the last one
        // sqrt(650 * 700); with three values, two stay above and one midpoint remains.
        let t = |i: usize| CuttingTest::new(format!("t{i}"), 2.0, 0.1e-3, 1e-3, 0.0).unwrap();
        let tests: Vec<CuttingTest> = (0..9).map(t).collect();
        let mut ctx = Context::of(&tests);
        ctx.bue_gate_c = Some((0..9).map(|i| 400.0 + 50.0 * i as f64).collect());
        let on = bue_onsets(&tests, &ctx);
        assert_eq!(on.len(), 6);
        assert!((on[5] - (650.0f64 * 700.0).sqrt()).abs() < 1e-9, "{on:?}");
        let tests3: Vec<CuttingTest> = (0..3).map(t).collect();
        let mut ctx3 = Context::of(&tests3);
        ctx3.bue_gate_c = Some(vec![400.0, 500.0, 600.0]);
        assert_eq!(bue_onsets(&tests3, &ctx3), vec![(400.0f64 * 500.0).sqrt()]);
    }

    #[test]
    fn bue_indicator_switches_at_onset() {
        // Logistic in ln V with width 0.1: at V = onset it is 1/2; at V = 2 onset it is 1/(1 + e^6.93).
        assert!((bue_indicator(80.0, 80.0) - 0.5).abs() < 1e-12);
        assert!(bue_indicator(160.0, 80.0) < 1e-3 && bue_indicator(40.0, 80.0) > 0.999);
    }
}
