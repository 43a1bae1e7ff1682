//! Unit tests of `physics`.

use super::*;

#[test]
fn grid_ends_at_the_upper_bound() {
    let g = sample_grid(20.0, 560.0, 100.0);
    assert_eq!(g.len(), 7);
    assert!((g[5] - 520.0).abs() < 1e-12 && (g[6] - 560.0).abs() < 1e-12);
    let h = sample_grid(20.0, 1220.0, 100.0);
    assert_eq!(h.len(), 13);
}

#[test]
fn eq17_mu_times_pressure_is_eq17_shear_stress() {
    // Independent check against the model's own Eq 17 implementation.
    let f = Friction::PressureDependentShear { m0: 0.9, beta_per_pa: 0.012e-6 };
    for p in [1e3, 1e6, 50e6, 400e6, 3e9] {
        let tau = f.shear_stress_pa(p, 144e6);
        let mu = eq17_mu(0.9, 0.012e-6, 144e6, p);
        assert!((mu * p - tau).abs() <= 1e-9 * tau, "{p}");
    }
    // P -> 0 limit m0 k beta: 0.9 * 144e6 * 0.012e-6 = 1.5552.
    assert!((eq17_mu(0.9, 0.012e-6, 144e6, 0.0) - 1.5552).abs() < 1e-12);
}

#[test]
fn interpolated_eq17_is_within_one_percent() {
    // Abaqus interpolates mu linearly between table pressures; the shear stress mu(P) P of the
    // interpolated table must stay within 1 % of Eq 17 everywhere on the standard grid, for the
    // paper's betas (0.0045/MPa steel, 0.012/MPa AA6082) and a steeper 0.02/MPa.
    let grid: Vec<f64> = crate::STANDARD_CONTACT_PRESSURES_MPA.iter().map(|p| p * 1e6).collect();
    let k = 300e6;
    for beta in [0.0045e-6, 0.012e-6, 0.02e-6] {
        let mut worst: f64 = 0.0;
        for w in grid.windows(2) {
            let (p0, p1) = (w[0], w[1]);
            let (m0, m1) = (eq17_mu(1.0, beta, k, p0), eq17_mu(1.0, beta, k, p1));
            for i in 1..20 {
                let p = p0 + (p1 - p0) * f64::from(i) / 20.0;
                let mu = m0 + (m1 - m0) * (p - p0) / (p1 - p0);
                let exact = eq17_mu(1.0, beta, k, p) * p;
                worst = worst.max((mu * p - exact).abs() / exact);
            }
        }
        assert!(worst <= 0.01, "beta {beta}: worst interpolation error {worst}");
        assert!(worst > 1e-4, "beta {beta}: the check must see the interpolation ({worst})");
    }
}

#[test]
fn local_k_falls_with_temperature_and_is_zero_at_melting() {
    // C38 Table 5 set; k(T) = sigma_JC(2, 1e4, T)/sqrt(3) (paper Eqs 14, 16, 17).
    let jc = JcParams::new(589e6, 145e6, 0.25, 0.069, 1.1, 1.0, 1460.0, 20.0).unwrap();
    let ks: Vec<f64> = [20.0, 400.0, 800.0, 1200.0].iter().map(|&t| local_shear_strength_pa(&jc, t)).collect();
    assert!(ks.windows(2).all(|w| w[1] < w[0]), "{ks:?}");
    // At 400 degC: (589 + 145 2^0.25)(1 + 0.069 ln 1e4)(1 - (380/1440)^1.1)/sqrt(3) = 552.93 MPa
    // (the table: 553 MPa).
    assert!((ks[1] / 1e6 - 552.93).abs() < 0.05, "{}", ks[1] / 1e6);
    assert!(local_shear_strength_pa(&jc, 1460.0).abs() < 1e-6);
}

#[test]
fn tabular_strains_interpolate_jc_within_one_percent() {
    // Linear interpolation of A + B eps^n between the standard strains (Abaqus *PLASTIC) against
    // the law itself, for the fixture JC sets: C38, 42CrMo4, AA6082 (paper Table 5) and AISI 1045
    // (Jaspers & Dautzenberg 2002), over eps in [0.001, 5].
    let s = crate::STANDARD_PLASTIC_STRAINS;
    for (a, b, n) in [(589.0, 145.0, 0.25), (530.0, 153.0, 0.25), (250.0, 61.0, 0.43), (553.1, 600.8, 0.234)] {
        let law = |e: f64| a + b * f64::powf(e, n);
        let mut worst: f64 = 0.0;
        for w in s.windows(2).filter(|w| w[0] >= 0.001) {
            for i in 1..200 {
                let e = w[0] + (w[1] - w[0]) * f64::from(i) / 200.0;
                let lin = law(w[0]) + (law(w[1]) - law(w[0])) * (e - w[0]) / (w[1] - w[0]);
                worst = worst.max((lin - law(e)).abs() / law(e));
            }
        }
        assert!(worst <= 0.01 && worst > 1e-4, "A {a}: worst {worst}");
    }
}

#[test]
fn names_with_commas_are_rejected() {
    assert!(check_name("C38").is_ok());
    assert!(check_name("C38,x").is_err());
    assert!(check_label("paper test 3").is_ok());
    assert!(check_label("a,b").is_err());
}
