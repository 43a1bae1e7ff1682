//! Criterion benchmark: one full diagnosis (baseline, screen, joint refits, nested
//! leave-one-condition-out) of a 3 x 3 feed x speed design with concealed edge ploughing
//! (design note Sec 4.4 Demo A: AISI 1045, h = 0.05/0.1/0.2 mm, V = 100/200/300 m/min, p_c = 15,
//! p_t = 35 N/mm). Target (issue 6): <= 2 s on the 2-core CI machine.
//!
//! Method and last numbers: `benches/README.md`.

use criterion::{criterion_group, criterion_main, Criterion};
use cutcal_diagnose::lite::{solve, Hooks, LiteConstants};
use cutcal_diagnose::simulator::JcBox;
use cutcal_diagnose::{diagnose, Config, LiteSimulator};
use cutcal_model::{CuttingTest, JcParams};

fn dataset() -> (Vec<CuttingTest>, LiteSimulator) {
    // Jaspers & Dautzenberg 2002 as the nominal set; the truth has A and C shifted.
    let jc = JcParams {
        a_pa: 553.1e6,
        b_pa: 600.8e6,
        n: 0.234,
        c: 0.0134,
        m: 1.0,
        eps0_per_s: 1.0,
        tm_c: 1460.0,
        tr_c: 25.0,
    };
    let k = LiteConstants {
        c0: 5.0,
        delta: 0.05,
        eta: 0.9,
        psi: 0.9,
        t_work_c: 25.0,
        rho_cp: 7862.0 * (420.0 + 0.504 * 25.0),
        conductivity: 52.61 - 0.0281 * 25.0,
    };
    let truth = JcParams { a_pa: 600e6, c: 0.016, ..jc };
    let hooks = Hooks { edge_fc_n_per_m: 15e3, edge_ft_n_per_m: 35e3, ..Hooks::NEUTRAL };
    let mut tests = Vec::new();
    let mut i = 0;
    for h in [0.05, 0.1, 0.2] {
        for v in [100.0, 200.0, 300.0] {
            i += 1;
            let t = CuttingTest::new(format!("{i}"), v / 60.0, h * 1e-3, 2e-3, 0.1).expect("valid test");
            let s = solve(&t, &truth, &k, &hooks).expect("lite solves");
            // Deterministic +-2 % pattern instead of random noise.
            let z = ((i * 7919) % 13) as f64 / 13.0 - 0.5;
            let t = t
                .with_forces(Some(s.fc_n_per_m * (1.0 + 0.04 * z)), Some(s.ft_n_per_m * (1.0 - 0.06 * z)))
                .and_then(|t| t.with_chip_thickness(Some(s.chip_m * (1.0 + 0.05 * z * z))))
                .expect("valid measurements");
            tests.push(t);
        }
    }
    (tests, LiteSimulator::with_constants(jc, k, &JcBox::wide(), true))
}

fn bench(c: &mut Criterion) {
    let (tests, sim) = dataset();
    let cfg = Config::standard("B");
    let mut g = c.benchmark_group("diagnose");
    g.sample_size(10);
    g.bench_function("d9_concealed_ploughing_nested_loco", |b| {
        b.iter(|| diagnose(&sim, &tests, &cfg).expect("diagnosis runs"))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
