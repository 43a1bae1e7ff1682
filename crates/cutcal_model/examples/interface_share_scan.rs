//! Where a smaller interface heat share still gives a cooler interface (`Physics::interface_heat_share`,
//! the tool's share of the frictional heat, Loewen & Shaw 1954, on Oxley 1989 Sec 4.3): over the
//! range of the property test `interface_heat_share_acts_as_psi` (`tests/it/oxley_props.rs`; AISI
//! 1045 of Lalwani et al. 2009 with the JC set of Jaspers & Dautzenberg 2002), prints the largest
//! share below 1, in steps of 0.005, whose interface is no cooler than Oxley's all-to-the-chip (or
//! whose solve fails), and the condition where it occurs.
//!
//! Run: `cargo run -p cutcal_model --release --example interface_share_scan`
#![allow(clippy::print_stdout)]

use cutcal_model::oxley::{self, CuttingConditions, OxleyOptions, Physics};
use cutcal_model::JcParams;

fn main() {
    let material = cutcal_model::reference::aisi1045_lalwani2009();
    let jc = JcParams::new(553.1e6, 600.8e6, 0.234, 0.0134, 1.0, 1.0, 1460.0, 25.0).expect("a valid JC set");
    // (largest share with no cooler interface, speed m/min, uncut thickness mm, rake deg)
    let mut worst = (0.0f64, 0.0, 0.0, 0.0);
    for speed_m_min in [100.0, 120.0, 150.0, 200.0, 300.0, 400.0] {
        for uncut_mm in [0.08, 0.1, 0.15, 0.2, 0.3] {
            for rake_deg in [-5.0, 0.0, 5.0, 8.0, 10.0] {
                let cond =
                    CuttingConditions::new(speed_m_min / 60.0, uncut_mm * 1e-3, 1e-3, f64::to_radians(rake_deg), 25.0)
                        .expect("valid conditions");
                let t_int = |share: f64| {
                    let physics = Physics { interface_heat_share: share, ..Physics::baseline() };
                    oxley::predict(&material, &jc, &cond, &OxleyOptions::wide(), &physics).map(|p| p.temperature_int_c)
                };
                let Ok(full) = t_int(1.0) else {
                    println!("{speed_m_min} m/min, {uncut_mm} mm, {rake_deg} deg: no solution with share 1");
                    continue;
                };
                let first_not_cooler = (1..=100)
                    .map(|k| 1.0 - 0.005 * f64::from(k))
                    .find(|&share| !matches!(t_int(share), Ok(t) if t < full))
                    .unwrap_or(0.0);
                if first_not_cooler > worst.0 {
                    worst = (first_not_cooler, speed_m_min, uncut_mm, rake_deg);
                }
            }
        }
    }
    println!(
        "largest share with an interface no cooler than share 1: {:.3} (at {} m/min, {} mm, {} deg)",
        worst.0, worst.1, worst.2, worst.3
    );
}
