//! Unit tests of `bootstrap`.

use super::*;

// C38 test 3 (paper Table 6): Fc = 224 N/mm, Ft = 186 N/mm, tc = 0.157 mm.
const NOMINAL: Measurement =
    Measurement { cutting_force_n_per_m: 224e3, feed_force_n_per_m: 186e3, chip_thickness_m: 0.157e-3 };

fn options(samples: usize) -> BootstrapOptions {
    BootstrapOptions {
        samples,
        seed: 7,
        uncertainty: RelativeUncertainty { force: 0.03, chip_thickness: 0.05 },
        choices: None,
    }
}

/// A stand-in identification with a known linear response: A = Fc/1000 MPa, B = Ft/1000 MPa,
/// n = 1000 tc (mm -> a number near 0.157), C and m fixed.
fn linear(s: &Sample) -> Result<JcParams, IdentError> {
    let m = &s.measurement;
    Ok(JcParams {
        a_pa: m.cutting_force_n_per_m * 1e3,
        b_pa: m.feed_force_n_per_m * 1e3,
        n: m.chip_thickness_m * 1e3,
        c: 0.069,
        m: 1.1,
        eps0_per_s: 1.0,
        tm_c: 1460.0,
        tr_c: 20.0,
    })
}

#[test]
fn spread_matches_the_stated_uncertainty() {
    let r = bootstrap(&NOMINAL, &options(4000), linear).unwrap();
    assert_eq!((r.succeeded, r.failed), (4000, 0));
    let a = &r.parameters[0];
    // A = 224 MPa x (1 + 0.03 z): mean 224, std 6.72; with 4000 samples the standard error of
    // the std is 6.72/sqrt(2 x 3999) = 0.075, so 5 % (0.34) is > 4 standard errors.
    assert!((a.mean - 224.0).abs() < 0.5, "{a:?}");
    assert!((a.std - 6.72).abs() < 0.34, "{a:?}");
    // Normal quantiles: 224 -/+ 1.96 x 6.72 = 210.8 / 237.2.
    assert!((a.q025 - 210.8).abs() < 1.0 && (a.q975 - 237.2).abs() < 1.0, "{a:?}");
    let n = &r.parameters[2];
    assert!((n.std / n.mean - 0.05).abs() < 0.0025, "{n:?}");
    // Independent draws: |rho(A, B)| small; C does not vary, so its correlations are None.
    assert!(r.correlation[0][1].unwrap().abs() < 0.06);
    assert!((r.correlation[0][0].unwrap() - 1.0).abs() < 1e-12);
    assert!(r.correlation[3].iter().all(Option::is_none));
}

#[test]
fn results_do_not_depend_on_the_thread_count() {
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| bootstrap(&NOMINAL, &options(257), linear).unwrap())
    };
    let (one, two, three) = (run(1), run(2), run(3));
    // Bit-identical, not approximately equal: the point is determinism.
    let bits = |r: &BootstrapReport| {
        r.parameters.iter().flat_map(|p| [p.mean, p.std, p.q025, p.q975]).map(f64::to_bits).collect::<Vec<_>>()
    };
    assert_eq!(bits(&one), bits(&two));
    assert_eq!(bits(&one), bits(&three));
    assert_ne!(bits(&one), bits(&pool_free_other_seed()));
}

fn pool_free_other_seed() -> BootstrapReport {
    bootstrap(&NOMINAL, &BootstrapOptions { seed: 8, ..options(257) }, linear).unwrap()
}

#[test]
fn choices_are_drawn_in_their_ranges_without_changing_the_measurements() {
    let c = UnstatedChoices::new([0.5, 2.0], 1.0).unwrap();
    let u = RelativeUncertainty { force: 0.03, chip_thickness: 0.05 };
    let (mut ln_h, mut r_sum) = (Vec::new(), 0.0);
    for i in 0..4000 {
        let s = sample(&NOMINAL, &u, Some(&c), 7, i);
        // The measurement is the one drawn without choices (same stream, drawn first).
        assert_eq!(s.measurement, perturbed(&NOMINAL, &u, 7, i));
        assert!((0.5..=2.0).contains(&s.h_factor) && (-1.0..=1.0).contains(&s.r_offset));
        ln_h.push(s.h_factor.ln());
        r_sum += s.r_offset;
    }
    // ln h uniform on [-ln 2, ln 2]: mean 0, sd ln2/sqrt 3 = 0.400; r uniform: mean 0.
    let (m, sd) = mean_std(&ln_h);
    assert!(m.abs() < 0.02 && (sd - 2f64.ln() / 3f64.sqrt()).abs() < 0.01, "{m} {sd}");
    assert!((r_sum / 4000.0).abs() < 0.03);
    let none = sample(&NOMINAL, &u, None, 7, 3);
    assert_eq!((none.h_factor, none.r_offset), (1.0, 0.0));
    assert!(UnstatedChoices::new([1.5, 2.0], 1.0).is_err());
    assert!(UnstatedChoices::new([0.5, 2.0], -1.0).is_err());
}

#[test]
fn failed_samples_are_counted_and_quoted() {
    let flaky = |s: &Sample| {
        let m = &s.measurement;
        if m.chip_thickness_m > 0.157e-3 {
            Err(IdentError::InvalidOptions("chip too thick".into()))
        } else {
            linear(s)
        }
    };
    let r = bootstrap(&NOMINAL, &options(400), flaky).unwrap();
    // About half of a symmetric perturbation lies above the nominal chip thickness.
    assert!(r.failed > 150 && r.failed < 250, "{}", r.failed);
    assert_eq!(r.succeeded + r.failed, 400);
    assert!(r.first_failure.as_deref().unwrap().contains("chip too thick"));
    let e = bootstrap(&NOMINAL, &options(10), |_| Err(IdentError::InvalidOptions("no".into()))).unwrap_err();
    assert!(e.to_string().contains("only 0 of 10"), "{e}");
}

#[test]
fn invalid_options_are_rejected() {
    assert!(bootstrap(&NOMINAL, &options(1), linear).is_err());
    let bad =
        BootstrapOptions { uncertainty: RelativeUncertainty { force: f64::NAN, chip_thickness: 0.05 }, ..options(10) };
    assert!(bootstrap(&NOMINAL, &bad, linear).unwrap_err().to_string().contains("force uncertainty"));
}

#[test]
fn quantile_interpolates_order_statistics() {
    // Type 7 on 1..=5: p = 0.1 -> h = 0.4 -> 1.4; p = 0.975 -> h = 3.9 -> 4.9.
    let x = [5.0, 1.0, 3.0, 2.0, 4.0];
    assert!((quantile(&x, 0.1) - 1.4).abs() < 1e-12);
    assert!((quantile(&x, 0.975) - 4.9).abs() < 1e-12);
}
