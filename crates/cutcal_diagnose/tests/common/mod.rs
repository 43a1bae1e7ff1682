//! Shared setup of the Mode A integration tests that read recordings through the full model:
//! the "external simulation" is cutcal's Oxley model on C38 thermal data (paper Table 3), the
//! shadow runs on generic steel (AISI 1045, Lalwani 2009), as in `mode_a.rs`.

#![allow(dead_code)]

use cutcal_diagnose::hooks::Hooks;
use cutcal_diagnose::simulator::oxley_with_hooks;
use cutcal_diagnose::{diagnose, Config, Prediction, ShadowSimulation};
use cutcal_model::oxley::OxleyOptions;
use cutcal_model::{CuttingTest, JcParams};

pub fn jaspers(room_c: f64) -> JcParams {
    JcParams::new(553.1e6, 600.8e6, 0.234, 0.0134, 1.0, 1.0, 1460.0, room_c).unwrap()
}

/// 3 feeds x 5 speeds at 0 deg rake, 2 mm wide; run order a fixed permutation (7 i mod 15) so that
/// it is not aligned with feed or speed.
pub fn design() -> Vec<CuttingTest> {
    let mut v = Vec::new();
    for (i, (h, s)) in
        [0.05, 0.1, 0.2].iter().flat_map(|h| [60.0, 100.0, 150.0, 220.0, 300.0].map(|s| (*h, s))).enumerate()
    {
        let mut t = CuttingTest::new(format!("{}", i + 1), s / 60.0, h * 1e-3, 2e-3, 0.0).unwrap();
        t.order = Some(((7 * i) % 15 + 1) as u32);
        v.push(t);
    }
    v
}

pub fn external(tests: &[CuttingTest], h: &dyn Fn(&CuttingTest) -> Hooks) -> Vec<Prediction> {
    let c38 = cutcal_model::reference::c38_table3();
    tests.iter().map(|t| oxley_with_hooks(&c38, &jaspers(20.0), t, &h(t), &OxleyOptions::wide()).unwrap()).collect()
}

/// Recordings from `rec` with both forces multiplied by `gain(test)` and a deterministic +-2 %
/// scatter (no random numbers: the test does not depend on a generator).
pub fn measured(tests: &[CuttingTest], rec: &[Prediction], gain: &dyn Fn(&CuttingTest) -> f64) -> Vec<CuttingTest> {
    tests
        .iter()
        .zip(rec)
        .enumerate()
        .map(|(i, (t, r))| {
            let z = ((i * 7919) % 13) as f64 / 13.0 - 0.5;
            let g = gain(t);
            t.clone()
                .with_forces(Some(r.fc_n_per_m * g * (1.0 + 0.04 * z)), Some(r.ft_n_per_m * g * (1.0 - 0.04 * z)))
                .and_then(|t| t.with_chip_thickness(Some(r.chip_m * (1.0 + 0.04 * z * z))))
                .unwrap()
        })
        .collect()
}

pub fn run(rec: &[CuttingTest], ext: &[Prediction]) -> cutcal_diagnose::Report {
    let sim = ShadowSimulation::build(&cutcal_model::reference::aisi1045_lalwani2009(), jaspers(25.0), rec, ext, true)
        .unwrap();
    diagnose(&sim, rec, &Config::standard("A")).unwrap()
}
