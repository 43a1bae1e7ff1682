//! Criterion benchmark (issue 10, "Speed"): one Mode A diagnosis of 15 conditions (3 feeds x 5
//! speeds), including the shadow fit of the external simulation, its signature tables and the
//! calibrated null (200 replicates, parallel). Target: <= 1 s on the 2-core CI machine.
//!
//! The "external simulation" is cutcal's Oxley model on C38 thermal data (paper Table 3) with the
//! Jaspers & Dautzenberg 2002 JC set; the recordings carry a 25 um edge (Waldorf et al. 1998) and a
//! deterministic +-2 % pattern. The shadow runs on generic steel (AISI 1045, Lalwani 2009).
//!
//! A second case runs the same data without a material file: every generic class's shadow is
//! built and fitted and the best one kept (`classes::best_shadow`), as the CLI does.
//!
//! Method and last numbers: `benches/README.md`.

use criterion::{criterion_group, criterion_main, Criterion};
use cutcal_diagnose::hooks::Hooks;
use cutcal_diagnose::simulator::oxley_with_hooks;
use cutcal_diagnose::{diagnose, Config, Prediction, ShadowSimulation};
use cutcal_model::oxley::OxleyOptions;
use cutcal_model::{CuttingTest, JcParams};

fn dataset() -> (Vec<CuttingTest>, Vec<Prediction>) {
    let jc = JcParams::new(553.1e6, 600.8e6, 0.234, 0.0134, 1.0, 1.0, 1460.0, 20.0).expect("valid JC");
    let mat = cutcal_model::reference::c38_table3();
    let o = OxleyOptions::wide();
    let edge = Hooks { edge_radius_m: 25e-6, ..Hooks::NEUTRAL };
    let (mut tests, mut ext) = (Vec::new(), Vec::new());
    let mut i = 0;
    for h in [0.05, 0.1, 0.2] {
        for v in [60.0, 100.0, 150.0, 220.0, 300.0] {
            i += 1;
            let t = CuttingTest::new(format!("{i}"), v / 60.0, h * 1e-3, 2e-3, 0.0).expect("valid test");
            let sim = oxley_with_hooks(&mat, &jc, &t, &Hooks::NEUTRAL, &o).expect("model solves");
            let rec = oxley_with_hooks(&mat, &jc, &t, &edge, &o).expect("model solves");
            let z = ((i * 7919) % 13) as f64 / 13.0 - 0.5;
            let t = t
                .with_forces(Some(rec.fc_n_per_m * (1.0 + 0.04 * z)), Some(rec.ft_n_per_m * (1.0 - 0.06 * z)))
                .and_then(|t| t.with_chip_thickness(Some(rec.chip_m * (1.0 + 0.05 * z * z))))
                .expect("valid measurements");
            tests.push(t);
            ext.push(sim);
        }
    }
    (tests, ext)
}

fn bench(c: &mut Criterion) {
    let (tests, ext) = dataset();
    let steel = cutcal_model::reference::aisi1045_lalwani2009();
    let jc = JcParams::new(553.1e6, 600.8e6, 0.234, 0.0134, 1.0, 1.0, 1460.0, 25.0).expect("valid JC");
    let cfg = Config::standard("A");
    let mut g = c.benchmark_group("diagnose");
    g.sample_size(10);
    g.bench_function("mode_a_15_conditions_shadow_and_calibrated_null", |b| {
        b.iter(|| {
            let sim = ShadowSimulation::build(&steel, jc, &tests, &ext, true).expect("shadow builds");
            diagnose(&sim, &tests, &cfg).expect("diagnosis runs")
        })
    });
    // The main Mode A case: no material file, so every generic class's shadow is built and fitted
    // and the best fitted one kept (`classes::best_shadow`) before the diagnosis.
    g.bench_function("mode_a_15_conditions_no_material_class_choice", |b| {
        b.iter(|| {
            let choice =
                cutcal_diagnose::classes::best_shadow(&tests, &ext, true, None).expect("a class's shadow builds");
            diagnose(&choice.shadow, &tests, &cfg).expect("diagnosis runs")
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
