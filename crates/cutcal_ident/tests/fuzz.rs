//! Property-based fuzzing of the DPZD identification: zones from random (mostly admissible)
//! shear-plane states, random bounds (sometimes inverted, NaN or infinite), random point and start
//! counts. Properties: no panic; an accepted identification is finite, inside its bounds and a
//! valid JC set.
//!
//! `CUTCAL_FUZZ_CASES` scales the case count (default: a bounded smoke run); see `docs/fuzzing.md`.
// Tests compare bit-identical results on purpose (determinism, warm against cold paths), print
// what they measure, and reject NaN with negated comparisons.
#![allow(clippy::float_cmp, clippy::print_stdout, clippy::print_stderr, clippy::neg_cmp_op_on_partial_ord)]

use cutcal_ident::{identify_from_zone, JcBounds, JcConstants, MultistartOptions};
use cutcal_model::dpzd::{self, DpzdConfig, DpzdVariant, ShearPlaneState};
use cutcal_model::Material;
use proptest::prelude::*;

fn config(smoke: u32) -> ProptestConfig {
    let cases = std::env::var("CUTCAL_FUZZ_CASES").ok().and_then(|s| s.parse().ok()).unwrap_or(smoke);
    ProptestConfig { cases, ..ProptestConfig::default() }
}

/// C38 of the paper's Table 3, in SI.
fn c38() -> Material {
    cutcal_model::reference::c38_table3()
}

/// A bound pair: usually sensible, sometimes inverted, negative, NaN or infinite.
fn pair(lo: f64, hi: f64) -> impl Strategy<Value = [f64; 2]> {
    prop_oneof![
        6 => (0.0f64..1.0, 0.0f64..1.0).prop_map(move |(a, b)| {
            let (x, y) = (lo + a * (hi - lo), lo + b * (hi - lo));
            [x.min(y), x.max(y)]
        }),
        1 => (any::<f64>(), any::<f64>()).prop_map(|(a, b)| [a, b]),
        1 => proptest::sample::select(vec![[f64::NAN, 1.0], [1.0, 0.5], [-1.0, 1.0], [0.0, f64::INFINITY], [0.3, 0.3]]),
    ]
}

proptest! {
    #![proptest_config(config(48))]

    #[test]
    fn identification_never_panics_and_respects_its_bounds(
        tau in 4.5e8f64..1.2e9, phi in 0.2f64..0.8, v in 0.5f64..8.0, enhanced in any::<bool>(),
        a in pair(1.0, 2000.0), b in pair(1.0, 2000.0), n in pair(0.0, 1.0), c in pair(0.0, 1.0), m in pair(0.0, 3.0),
        points in 0usize..60, starts in 0usize..4, seed in any::<u64>(),
    ) {
        let variant = if enhanced {
            DpzdVariant::Enhanced { tolerance_c: 1e-6, max_iterations: 50 }
        } else {
            DpzdVariant::Original { rho_cp_j_per_m3_k: 3.5325e6 }
        };
        let cfg = DpzdConfig::new(1e-4, 4.0, variant).expect("paper Sec 4.2 settings");
        let state = ShearPlaneState { speed_m_per_s: v, rake_rad: 0.0, shear_angle_rad: phi, tau_max_pa: tau };
        let Ok(zone) = dpzd::solve(&c38(), &state, &cfg) else { return Ok(()) };
        let bounds = JcBounds { a_mpa: a, b_mpa: b, n, c, m };
        let constants = JcConstants { eps0_per_s: 1.0, tm_c: 1460.0, tr_c: 20.0 };
        let options = MultistartOptions::new(starts, seed);
        if let Ok(id) = identify_from_zone(&zone, points, &bounds, constants, &options) {
            prop_assert!(id.jc.validate().is_ok(), "{:?}", id.jc);
            prop_assert!(id.objective_mpa.is_finite() && id.rms_mpa.is_finite());
            // Compared in the units the identification stores (Pa): MPa -> Pa -> MPa does not round-trip.
            let got = [id.jc.a_pa, id.jc.b_pa, id.jc.n, id.jc.c, id.jc.m];
            let scale = [1e6, 1e6, 1.0, 1.0, 1.0];
            for ((v, [lo, hi]), k) in got.iter().zip([a, b, n, c, m]).zip(scale) {
                prop_assert!(*v >= lo * k && *v <= hi * k, "{} outside [{}, {}]", v, lo * k, hi * k);
            }
            prop_assert!(points >= 6 && starts >= 1);
        }
    }
}
