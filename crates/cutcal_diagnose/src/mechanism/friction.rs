//! The tool-chip friction law of the friction mechanism (design note M4, M5): the shear factor
//! `m_f0 (V / V_ref)^(-p_v)` and its second form, the hybrid Coulomb-Tresca cap
//! (`screen::coulomb_form` refits both and keeps the better).

/// Speed-dependent interface friction factor `m_f0 (V / V_ref)^(-p_v)` (design note M5, the power
/// law in V; Rech, Claudin & D'Eramo 2009 measured friction falling with sliding speed).
#[must_use]
pub fn friction_factor(m_f0: f64, p_v: f64, speed_m_min: f64, v_ref_m_min: f64) -> f64 {
    m_f0 * (speed_m_min / v_ref_m_min).powf(-p_v)
}

/// The interface friction factor of a test whose baseline friction load is `load` (its apparent
/// coefficient `k_chip / sigma_N` over the dataset's largest, `Context::friction_load`), with the
/// Coulomb share `w_c` (the mechanism uses 0 or 1 as `Context::friction_coulomb` is false or true):
/// `min(1, m (1 / load)^w_c)`, `m` from [`friction_factor`].
///
/// At `w_c = 0` the factor is the constant (or speed-dependent) `m` of the shear-factor law. At
/// `w_c = 1` it is the hybrid Coulomb-Tresca law `tau_int = min(mu sigma_N, k_chip)` (Zorev 1963;
/// the law of DEFORM and Abaqus, Oezel 2006, Int. J. Mach. Tools Manuf. 46, 518) with `mu = m
/// mu_max`: the interface slides where the baseline needs more than `mu` to stick (the test of
/// largest load, a cool chip on a hard primary zone) and sticks, unchanged, where it needs less.
/// Taken at the baseline's stresses (the first step of the fixed point; the cap lowers the chip's
/// temperature and so raises `k_chip` a little, which the twenty-seventh session measured as a
/// narrower range of factors when solved: 0.82-1 against 0.57-1). At `m = 1` the factor is 1 for every `w_c`.
#[must_use]
pub fn hybrid_friction_factor(m: f64, load: f64, w_c: f64) -> f64 {
    (m * load.clamp(1e-3, 1.0).powf(-w_c.clamp(0.0, 1.0))).min(1.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hooks::Hooks;
    use crate::mechanism::{set_hooks, Context, MechanismId};
    use crate::simulator::Simulator;
    use cutcal_model::CuttingTest;

    #[test]
    fn friction_factor_falls_with_speed_about_the_reference() {
        // m_f0 (V/V_ref)^(-p_v): equal to m_f0 at V_ref, 2^(-0.2) = 0.8706 of it at twice V_ref,
        // constant when p_v = 0; the context's V_ref is the geometric mean speed (80, 320 -> 160).
        assert!((friction_factor(0.7, 0.2, 150.0, 150.0) - 0.7).abs() < 1e-12);
        assert!((friction_factor(0.7, 0.2, 300.0, 150.0) - 0.7 * 0.870_550_563_3).abs() < 1e-9);
        assert!((friction_factor(0.7, 0.0, 37.0, 150.0) - 0.7).abs() < 1e-12);
        let tests = [
            CuttingTest::new("a", 80.0 / 60.0, 0.1e-3, 1e-3, 0.0).unwrap(),
            CuttingTest::new("b", 320.0 / 60.0, 0.1e-3, 1e-3, 0.0).unwrap(),
        ];
        assert!((Context::of(&tests).friction_v_ref_m_min - 160.0).abs() < 1e-9);
    }

    #[test]
    fn speed_exponent_moves_the_oxley_model_in_the_m5_direction() {
        // Note Sec 2.3, M5: with p_v > 0 the feed force falls with ln V relative to constant m_f.
        let m = cutcal_model::reference::aisi1045_lalwani2009();
        let jc = crate::simulator::tests::jaspers();
        let tests = [
            CuttingTest::new("lo", 100.0 / 60.0, 0.1e-3, 1e-3, 0.0).unwrap(),
            CuttingTest::new("hi", 400.0 / 60.0, 0.1e-3, 1e-3, 0.0).unwrap(),
        ];
        let ctx = Context::of(&tests);
        let sim = crate::simulator::OxleySimulator::new(&m, jc, &crate::simulator::JcBox::wide(), false);
        let ratio = |p_v: f64| {
            let mut hooks = [Hooks::NEUTRAL; 2];
            set_hooks(MechanismId::ToolChipFriction, &[0.7, p_v], &tests, &ctx, &sim, &mut hooks);
            let r = sim.simulate(&tests, &[], &hooks).unwrap();
            r[1].ft_n_per_m / r[0].ft_n_per_m
        };
        assert!(ratio(0.3) < 0.97 * ratio(0.0), "{} vs {}", ratio(0.3), ratio(0.0));
    }

    #[test]
    fn the_coulomb_share_caps_friction_where_the_load_is_high_and_never_beyond_sticking() {
        // min(1, m load^(-w_c)), by hand: with m = 0.6, w_c = 1 the largest load (1) keeps 0.6,
        // a load of 0.8 gives 0.6 / 0.8 = 0.75, and one of 0.5 would give 1.2, so it sticks (1).
        assert!((hybrid_friction_factor(0.6, 1.0, 1.0) - 0.6).abs() < 1e-12);
        assert!((hybrid_friction_factor(0.6, 0.8, 1.0) - 0.75).abs() < 1e-12);
        assert!((hybrid_friction_factor(0.6, 0.5, 1.0) - 1.0).abs() < 1e-12);
        // w_c = 1/2 takes the square root of the load: 0.6 / sqrt(0.64) = 0.75.
        assert!((hybrid_friction_factor(0.6, 0.64, 0.5) - 0.75).abs() < 1e-12);
        // w_c = 0 is the shear-factor law, and at m = 1 the law is off at any share.
        assert!((hybrid_friction_factor(0.6, 0.3, 0.0) - 0.6).abs() < 1e-12);
        for w in [0.0, 0.3, 1.0] {
            assert!((hybrid_friction_factor(1.0, 0.3, w) - 1.0).abs() < 1e-12);
        }
    }
}
