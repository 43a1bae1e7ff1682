//! Benchmark: one extended Oxley prediction (Lalwani et al. 2009, AISI 1045 case 1), cold start.
use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use cutcal_model::oxley::{self, CuttingConditions, OxleyOptions, Physics};
use cutcal_model::{JcParams, Material, TempPolynomial, ThermalProperties};

fn aisi1045() -> Material {
    // Lalwani et al. 2009: rho 7862 kg/m3, Cp = 420 + 0.504 T, K = 52.61 - 0.0281 T.
    let rho = TempPolynomial::constant(7862.0);
    Material {
        name: "AISI1045".into(),
        thermal: ThermalProperties {
            rho_cp: rho.product(&TempPolynomial::new(vec![420.0, 0.504]).unwrap()),
            density: rho,
            conductivity: TempPolynomial::new(vec![52.61, -0.0281]).unwrap(),
            valid_from_c: 0.0,
            valid_to_c: 1400.0,
        },
        yield_strength: None,
        melting_c: 1460.0,
        room_c: 25.0,
        elastic: None,
    }
}

fn bench(c: &mut Criterion) {
    let m = aisi1045();
    // Jaspers & Dautzenberg 2002.
    let jc = JcParams::new(553.1e6, 600.8e6, 0.234, 0.0134, 1.0, 1.0, 1460.0, 25.0).unwrap();
    let cond = CuttingConditions::new(200.0 / 60.0, 0.15e-3, 1.6e-3, (-7f64).to_radians(), 25.0).unwrap();
    let opts = OxleyOptions::wide();
    let phys = Physics::baseline();
    c.bench_function("oxley_predict_aisi1045_case1", |b| {
        b.iter(|| oxley::predict(black_box(&m), black_box(&jc), black_box(&cond), &opts, &phys).unwrap())
    });
    let start = oxley::predict(&m, &jc, &cond, &opts, &phys).unwrap();
    c.bench_function("oxley_predict_aisi1045_case1_warm", |b| {
        b.iter(|| oxley::predict_from(black_box(&m), black_box(&jc), &cond, &opts, &phys, Some(&start)).unwrap())
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
