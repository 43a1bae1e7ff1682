//! Synthetic recordings with known truth: window, mean, sd, drift and oscillation flags.
//!
//! The truth is the generator's input (`SyntheticSpec`): levels, noise sd, ramps, drift and the
//! oscillation are set, never fitted. Tolerances are those of issue 13 (mean 0.5 %, sd 10 %).
// Tests compare bit-identical results on purpose (determinism, warm against cold paths), print
// what they measure, and reject NaN with negated comparisons.
#![allow(clippy::float_cmp, clippy::print_stdout, clippy::print_stderr, clippy::neg_cmp_op_on_partial_ord)]

use cutcal_signal::synthetic::SyntheticSpec;
use cutcal_signal::{analyse, Analysis, AnalysisConfig, Reduced, DEFAULT_MAX_BLOCKS};
use proptest::prelude::*;

fn run(spec: &SyntheticSpec) -> Analysis {
    let r = Reduced::from_samples(3, DEFAULT_MAX_BLOCKS, spec.samples()).unwrap();
    analyse(&r, &AnalysisConfig::default(), None).unwrap()
}

/// Mean of the truth over the detected window (it differs from the level when there is a drift).
fn true_mean(spec: &SyntheticSpec, c: usize, a: &Analysis) -> f64 {
    let n = 20_000;
    (0..n).map(|i| spec.truth(c, a.t0_s + (a.t1_s - a.t0_s) * (i as f64 + 0.5) / n as f64)).sum::<f64>() / n as f64
}

fn check_window_and_moments(spec: &SyntheticSpec, a: &Analysis) {
    check_window_and_moments_tol(spec, a, 0.0);
}

/// `se_factor > 0`: with strongly correlated noise the sampling error of a 1.5 s cut can exceed
/// 0.5 %; the mean must then lie within `se_factor` reported standard errors of the truth (which
/// also checks that the standard error is honest).
fn check_window_and_moments_tol(spec: &SyntheticSpec, a: &Analysis, se_factor: f64) {
    let (s0, s1) = spec.steady();
    assert!(a.t0_s >= s0 && a.t1_s <= s1, "window {:.4}..{:.4} not inside steady {s0}..{s1}", a.t0_s, a.t1_s);
    assert!(a.t1_s - a.t0_s > 0.8 * (s1 - s0), "window {:.4}..{:.4} keeps < 80 % of the cut", a.t0_s, a.t1_s);
    for c in 0..3 {
        let m = true_mean(spec, c, a);
        let got = a.channels[c].mean;
        let tol = (0.005 * m).max(se_factor * a.channels[c].se);
        assert!((got - m).abs() <= tol, "channel {c}: mean {got} vs truth {m} (se {})", a.channels[c].se);
    }
}

#[test]
fn plain_cut_mean_sd_and_no_flags() {
    let spec = SyntheticSpec::plain(11);
    let a = run(&spec);
    check_window_and_moments(&spec, &a);
    for c in 0..3 {
        let sd = a.channels[c].sd;
        assert!((sd - spec.noise_sd_n[c]).abs() <= 0.10 * spec.noise_sd_n[c], "channel {c}: sd {sd}");
        // White noise: the standard error is sd / sqrt(n) within the estimator's spread.
        let iid = sd / (a.samples_used as f64).sqrt();
        assert!(a.channels[c].se < 1.6 * iid, "channel {c}: se {} vs iid {iid}", a.channels[c].se);
    }
    assert!(!a.possible_tool_wear && !a.possible_built_up_edge, "{a:?}");
}

#[test]
fn correlated_noise_inflates_the_standard_error() {
    // AR(1) phi = 0.9: tau = (1 + phi) / (1 - phi) = 19, so se = sd * sqrt(19 / n).
    let spec = SyntheticSpec { noise_phi: 0.9, ..SyntheticSpec::plain(3) };
    let a = run(&spec);
    check_window_and_moments(&spec, &a);
    let ch = a.channels[0];
    let expect = ch.sd * (19.0 / a.samples_used as f64).sqrt();
    assert!((ch.se / expect - 1.0).abs() < 0.35, "se {} vs AR(1) value {expect}", ch.se);
    assert!((ch.sd - 10.0).abs() <= 1.0, "sd {}", ch.sd);
    assert!(!a.possible_tool_wear && !a.possible_built_up_edge);
}

#[test]
fn drift_is_flagged() {
    let spec = SyntheticSpec { drift_relative: 0.08, ..SyntheticSpec::plain(5) };
    let a = run(&spec);
    check_window_and_moments(&spec, &a);
    assert!(a.possible_tool_wear, "{:?}", a.channels[0]);
    // Slope truth: 8 % of 500 N over 1.45 s.
    let slope = 0.08 * 500.0 / 1.45;
    assert!((a.channels[0].drift_per_s / slope - 1.0).abs() < 0.1, "slope {}", a.channels[0].drift_per_s);
    assert!(!a.possible_built_up_edge);
}

#[test]
fn bue_oscillation_is_flagged_with_its_frequency_and_amplitude() {
    let spec = SyntheticSpec { oscillation: Some((45.0, 0.08)), ..SyntheticSpec::plain(9) };
    let a = run(&spec);
    check_window_and_moments(&spec, &a);
    let ch = a.channels[0];
    assert!(a.possible_built_up_edge, "{ch:?}");
    assert!((ch.oscillation_hz.unwrap() - 45.0).abs() < 1.0, "{ch:?}");
    assert!((ch.oscillation_amplitude.unwrap() / 40.0 - 1.0).abs() < 0.1, "{ch:?}");
    assert!(!a.possible_tool_wear, "{ch:?}");
    // sd of noise + sinusoid: sqrt(10^2 + 40^2 / 2).
    let sd = (100.0f64 + 800.0).sqrt();
    assert!((ch.sd / sd - 1.0).abs() < 0.1, "{ch:?}");
}

#[test]
fn dropout_is_excluded() {
    let spec = SyntheticSpec { dropout: Some((0.9, 0.01)), ..SyntheticSpec::plain(13) };
    let a = run(&spec);
    check_window_and_moments(&spec, &a);
    assert_eq!(a.samples_dropped, 100);
    assert!((a.channels[0].sd - 10.0).abs() <= 1.0);
    assert!(!a.possible_tool_wear && !a.possible_built_up_edge);
}

#[test]
fn slow_ramps_and_a_long_idle_record() {
    let spec = SyntheticSpec {
        duration_s: 6.0,
        entry_s: 1.5,
        ramp_s: 0.3,
        exit_s: 4.0,
        rate_hz: 2_000.0,
        ..SyntheticSpec::plain(21)
    };
    let a = run(&spec);
    check_window_and_moments(&spec, &a);
}

#[test]
fn high_rate_long_record_is_decimated() {
    // 100 kHz, 3 s: more samples than blocks, so the block length grows.
    let spec = SyntheticSpec { rate_hz: 100_000.0, duration_s: 3.0, exit_s: 2.6, ..SyntheticSpec::plain(4) };
    let a = run(&spec);
    assert!(a.block_len > 1);
    check_window_and_moments(&spec, &a);
}

#[test]
fn given_window_is_used() {
    let spec = SyntheticSpec::plain(2);
    let r = Reduced::from_samples(3, DEFAULT_MAX_BLOCKS, spec.samples()).unwrap();
    let a = analyse(&r, &AnalysisConfig::default(), Some((0.5, 1.0))).unwrap();
    assert!(a.window_given);
    assert!((a.t0_s - 0.5).abs() < 1e-3 && (a.t1_s - 1.0).abs() < 1e-3, "{} {}", a.t0_s, a.t1_s);
    assert!((a.channels[0].mean / 500.0 - 1.0).abs() < 0.005);
}

#[test]
fn all_zero_signal_is_no_cut() {
    let r = Reduced::from_samples(1, 64, (0..1000).map(|i| (i as f64 * 1e-3, [0.0]))).unwrap();
    assert!(analyse(&r, &AnalysisConfig::default(), None).is_err());
}

/// False alarms are a rate, not an impossibility: the drift flag tests |z| > 3.29, a two-sided level
/// of 0.001 (and a change above 2 % of the mean), so noise alone may raise it about once in a
/// thousand signals, and less where the change stays under 2 %. Over 800 noise-only signals (white
/// and AR(1) noise, phi 0-0.95, sd 0.5-6 % of the mean, fixed seeds) each flag is raised at most 4
/// times: with the level 0.001, Binomial(800, 0.001) exceeds 4 with probability 0.0014, while a
/// standard error 30 % too small (3.29 reached at a true z of 2.3, p 0.021) would let the z test
/// pass about 17 times before the 2 % condition. The built-up-edge flag has no stated level; it is held to the same rate. Measured
/// once over 4000 other seeds of the same grid: 1 drift flag, and 3 built-up-edge flags, all at
/// phi 0.95 with 6 % noise (3 of 250 there: a strongly red spectrum can stand a low line 8x above
/// the band median).
#[test]
fn noise_alone_raises_a_flag_no_more_often_than_the_drift_level() {
    let (mut wear, mut bue) = (Vec::new(), Vec::new());
    for i in 0..800u64 {
        let phi = [0.0, 0.5, 0.8, 0.95][(i % 4) as usize];
        let rel_sd = [0.005, 0.02, 0.04, 0.06][((i / 4) % 4) as usize];
        let spec = SyntheticSpec {
            noise_phi: phi,
            noise_sd_n: [500.0 * rel_sd, 300.0 * rel_sd, 50.0 * rel_sd],
            rate_hz: 5_000.0,
            ..SyntheticSpec::plain(i)
        };
        let a = run(&spec);
        if a.possible_tool_wear {
            wear.push((i, phi, rel_sd, a.channels[0].drift_z));
        }
        if a.possible_built_up_edge {
            bue.push((i, phi, rel_sd, a.channels[0].oscillation_prominence));
        }
    }
    println!("noise only, 800 signals: drift flags {wear:?}; built-up-edge flags {bue:?}");
    assert!(wear.len() <= 4, "drift flags on noise alone: {wear:?}");
    assert!(bue.len() <= 4, "built-up-edge flags on noise alone: {bue:?}");
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, ..ProptestConfig::default() })]

    /// Noise only (white or correlated): the window and the moments are right. How often noise
    /// alone raises a flag is a rate, checked by `noise_alone_raises_a_flag_no_more_often_than_the_drift_level`:
    /// this property once claimed "never", and a 1000-seed audit (forty-third session) found a
    /// drift flag on AR(1) noise (audit seed 919: the signal's seed 2461, phi 0.77, sd 4.7 %,
    /// z 3.84, 2.1 % across the window).
    #[test]
    fn noise_alone_keeps_the_window_and_the_moments(seed in 0u64..10_000, phi in 0.0f64..0.95, rel_sd in 0.005f64..0.06) {
        let spec = SyntheticSpec { noise_phi: phi, noise_sd_n: [500.0 * rel_sd, 300.0 * rel_sd, 50.0 * rel_sd], rate_hz: 5_000.0, ..SyntheticSpec::plain(seed) };
        let a = run(&spec);
        check_window_and_moments_tol(&spec, &a, 4.0);
    }

    /// Detection: a drift of 5-15 % or an oscillation of 5-15 % at 20-200 Hz is always flagged,
    /// and only its own flag is raised.
    #[test]
    fn flags_when_present(seed in 0u64..10_000, drift in 0.05f64..0.15, f in 20.0f64..200.0, amp in 0.05f64..0.15, which in 0u8..2) {
        let base = SyntheticSpec { rate_hz: 5_000.0, ..SyntheticSpec::plain(seed) };
        if which == 0 {
            let a = run(&SyntheticSpec { drift_relative: drift, ..base });
            prop_assert!(a.possible_tool_wear && !a.possible_built_up_edge, "{:?}", a.channels[0]);
        } else {
            let a = run(&SyntheticSpec { oscillation: Some((f, amp)), ..base });
            prop_assert!(a.possible_built_up_edge && !a.possible_tool_wear, "{:?}", a.channels[0]);
            prop_assert!((a.channels[0].oscillation_hz.unwrap() - f).abs() < 1.5);
        }
    }
}
