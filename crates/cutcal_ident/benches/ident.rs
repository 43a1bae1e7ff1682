//! Benchmarks: one 50-start enhanced-DPZD identification of C38 test 3 (paper Table 4).
use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use cutcal_ident::{identify_from_zone, JcBounds, JcConstants, MultistartOptions};
use cutcal_model::dpzd::{self, DpzdConfig, DpzdVariant, ShearPlaneState};
use cutcal_model::{Material, TempPolynomial, ThermalProperties};

fn c38() -> Material {
    // Table 3 (paper), C38, SI.
    let rho = TempPolynomial::new(vec![7.866, -8.465e-4, 1.091e-6, -5.961e-10]).unwrap().scaled(1e3);
    let cp = TempPolynomial::new(vec![0.2306, 0.0025, -3.653e-6, 1.707e-9]).unwrap().scaled(1e3);
    Material {
        name: "C38".into(),
        thermal: ThermalProperties {
            rho_cp: rho.product(&cp),
            density: rho,
            conductivity: TempPolynomial::new(vec![45.1088, -0.0321, 1.645e-5]).unwrap(),
            valid_from_c: 20.0,
            valid_to_c: 1200.0,
        },
        yield_strength: Some(TempPolynomial::new(vec![773.007, -1.630, 0.0038, -3.001e-6]).unwrap().scaled(1e6)),
        melting_c: 1460.0,
        room_c: 20.0,
        elastic: None,
    }
}

fn bench(c: &mut Criterion) {
    let m = c38();
    let state = ShearPlaneState {
        speed_m_per_s: 4.0,
        rake_rad: 0.0,
        shear_angle_rad: (0.075f64 / 0.157).atan(),
        tau_max_pa: 700.9e6,
    };
    let cfg = DpzdConfig::new(1e-4, 4.0, DpzdVariant::Enhanced { tolerance_c: 1e-6, max_iterations: 50 }).unwrap();
    let z = dpzd::solve(&m, &state, &cfg).unwrap();
    let bounds = JcBounds { a_mpa: [1.0, 2000.0], b_mpa: [1.0, 2000.0], n: [0.0, 0.25], c: [1e-4, 1.0], m: [0.9, 1.1] };
    let consts = JcConstants { eps0_per_s: 1.0, tm_c: 1460.0, tr_c: 20.0 };
    let opts = MultistartOptions::new(50, 1);
    c.bench_function("identify_enhanced_c38_test3_50_starts", |b| {
        b.iter(|| identify_from_zone(black_box(&z), 51, &bounds, consts, &opts).unwrap())
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
